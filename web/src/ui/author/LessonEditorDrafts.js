// Drafts of lessons kept in this browser until they are saved: a page closed by mistake, or a
// sign-in that ran out before the save, loses no edits. A draft is kept with the ETag of the
// version it was made on, so that saving it over a newer version is a 412 like any stale save.

import { draftOf } from './LessonEditorModel.js';

/** The localStorage key under which drafts are kept (`.ID`, or `.new` for a lesson not saved yet). */
export const DRAFT_KEY = 'glasshead.lessonDraft';

/** The key of lesson `id`'s draft (null: a new lesson). */
export function draftKey( id ) {

	return `${ DRAFT_KEY }.${ id ?? 'new' }`;

}

function storage( win ) {

	try {

		return win?.localStorage ?? null;

	} catch {

		return null; // storage turned off: drafts live on the page only

	}

}

/** Keep `draft` of lesson `id`, made on the version `etag`. */
export function keepDraft( win, id, draft, etag ) {

	try {

		storage( win )?.setItem( draftKey( id ), JSON.stringify( { draft, etag } ) );

	} catch {
		// Full: the draft stays on the page only.
	}

}

/** Forget lesson `id`'s draft (it was saved, or dropped on purpose). */
export function forgetDraft( win, id ) {

	storage( win )?.removeItem( draftKey( id ) );

}

/** Lesson `id`'s kept draft, { draft, etag }, or null (none, or unreadable). */
export function keptDraft( win, id ) {

	try {

		const kept = JSON.parse( storage( win )?.getItem( draftKey( id ) ) ?? 'null' );
		return Array.isArray( kept?.draft?.items ) && kept.draft.items.length ? { draft: draftOf( kept.draft ), etag: kept.etag ?? null } : null;

	} catch {

		return null;

	}

}
