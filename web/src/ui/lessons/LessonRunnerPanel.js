// The lesson runner's side panel, for the teacher and hidden in presentation mode: give the lesson
// to one of their classes (GET /classes, POST /assignments) and see that class's practice of it
// (GET /children?class_id=, GET /practice?child_id=&lesson_id= for each child: newest first),
// each record with the child's picture and name, the item, how it went and when. Classes shared
// with the signed-in teacher or clinician are listed with their own; the class's owner shares it
// from here (LessonRunnerStaff.js).

import { h } from '../shared/dom.js';
import { picture, RATINGS } from '../shared/ChildPracticePictures.js';
import { targetLabel } from './LessonRunnerItems.js';
import { LessonRunnerJoin } from './LessonRunnerJoin.js';
import { LessonRunnerRoster } from './LessonRunnerRoster.js';
import { LessonRunnerStaff } from './LessonRunnerStaff.js';
import { isForbidden } from '../shared/signIn.js';

/** Records listed per child at most (the newest). */
const PER_CHILD = 50;

/**
 * The practice table's rows, newest first: { child, item, target, rating, replays, when } from
 * the records, the children ({ id, display_name, avatar }) and the lesson's items.
 */
export function practiceRows( records, children, items ) {

	const byId = new Map( children.map( ( child ) => [ child.id, child ] ) );
	return records
		.filter( ( record ) => byId.has( record.child_id ) )
		.sort( ( a, b ) => Date.parse( b.practised_at ) - Date.parse( a.practised_at ) || b.id - a.id )
		.map( ( record ) => ( {
			id: record.id,
			child: byId.get( record.child_id ),
			item: record.item_index,
			target: items[ record.item_index ] ? targetLabel( items[ record.item_index ] ) : `item ${ record.item_index + 1 }`,
			rating: RATINGS.find( ( r ) => r.rating === record.rating ) ?? null,
			ratedBy: record.rated_by,
			replays: record.replays,
			when: record.practised_at,
		} ) );

}

/** A time as the teacher reads it: today's as hours and minutes, an older one with its date. */
export function shortTime( iso, now = new Date() ) {

	const date = new Date( iso );
	const time = date.toLocaleTimeString( [], { hour: '2-digit', minute: '2-digit' } );
	return date.toDateString() === now.toDateString() ? time : `${ date.toLocaleDateString() } ${ time }`;

}

export class LessonRunnerPanel {

	/** @param {{ api: object }} options the page's API client */
	constructor( { api } ) {

		this.api = api;
		this.lesson = null;
		this.classes = [];
		this.rows = [];
		this.assigned = [];
		this.loads = 0;
		this.classSelect = h( 'select', { id: 'lr-class', className: 'lr-select', 'aria-label': 'Class', onChange: () => this.refresh() } );
		this.assignButton = h( 'button', { type: 'button', className: 'lr-assign', onClick: () => this.assign() }, 'Assign to this class' );
		this.assignedNote = h( 'p', { className: 'lr-note', role: 'status', 'aria-live': 'polite' } );
		this.join = new LessonRunnerJoin( { api } );
		this.childrenNote = h( 'p', { className: 'lr-note lr-children' } );
		this.roster = new LessonRunnerRoster( { api, classId: () => this.classId, onClass: ( made ) => this.loadClasses( made.id ), onChild: () => this.refresh() } );
		this.sharing = new LessonRunnerStaff( { api } );
		this.refreshButton = h( 'button', { type: 'button', onClick: () => this.refresh() }, 'Refresh' );
		this.table = h( 'ul', { className: 'lr-records', 'aria-label': 'Practice records' } );
		this.error = h( 'p', { className: 'error', role: 'alert', hidden: '' } );
		this.classLabel = h( 'label', { className: 'field-label', for: 'lr-class' }, 'Class' );
		this.recordsHead = h( 'div', { className: 'lr-records-head' }, h( 'h2', { className: 'lr-heading' }, 'Practice' ), this.refreshButton );
		this.element = h( 'aside', { className: 'lr-panel', 'aria-label': 'Class and practice' },
			this.classLabel, this.classSelect, this.assignButton, this.assignedNote, this.join.element, this.childrenNote, this.roster.element,
			this.sharing.element, this.recordsHead, this.table, this.error );

	}

	/** Show the panel for `lesson` ({ id, title, items }): the teacher's classes, then the practice. */
	async setLesson( lesson ) {

		this.lesson = lesson;
		await this.loadClasses();

	}

	/** The teacher's classes in the chooser (`chosen` chosen, else the one chosen before), then the practice. */
	async loadClasses( chosen = this.classSelect.value ) {

		try {

			this.classes = ( await this.api.get( 'classes?limit=100' ) ).classes ?? [];

		} catch ( error ) {

			this.classes = [];
			if ( isForbidden( error ) ) {

				// An author: lessons to run, but no classes to give them to.
				for ( const element of [ this.classLabel, this.classSelect, this.assignButton, this.roster.element, this.sharing.element, this.recordsHead, this.table ] ) element.hidden = true;
				this.assignedNote.textContent = 'Teachers, clinicians and admins give lessons to their classes here.';
				return;

			}

			this.showError( `Your classes could not be loaded: ${ error.message }` );

		}

		this.classSelect.replaceChildren( ...this.classes.map( ( c ) => h( 'option', { value: String( c.id ) }, c.name ) ) );
		if ( this.classes.some( ( c ) => String( c.id ) === String( chosen ) ) ) this.classSelect.value = String( chosen );
		const none = this.classes.length === 0;
		this.classSelect.disabled = none;
		this.assignButton.disabled = none;
		if ( none ) this.assignedNote.textContent = 'You have no classes yet: make one below.';
		this.roster.load( ! none );
		await this.refresh();

	}

	get classId() {

		return this.classSelect.value ? Number( this.classSelect.value ) : null;

	}

	/** Whether the chosen class has the lesson, and its children's practice of it. */
	async refresh() {

		const lesson = this.lesson;
		const classId = this.classId;
		const load = ++ this.loads;
		if ( classId !== this.sharing.classId ) this.sharing.load( classId ); // its own errors, its own line
		if ( ! lesson || classId === null ) {

			this.join.show( null );
			this.childrenNote.textContent = '';
			return this.show( [] );

		}

		this.showError( '' );
		try {

			const [ assignments, children ] = await Promise.all( [
				this.api.get( `assignments?lesson_id=${ lesson.id }&class_id=${ classId }` ),
				this.api.get( `children?class_id=${ classId }&limit=100` ),
			] );
			const kids = children.children ?? [];
			const lists = await Promise.all( kids.map( ( child ) => this.api.get( `practice?child_id=${ child.id }&lesson_id=${ lesson.id }&limit=${ PER_CHILD }` ) ) );
			if ( load !== this.loads ) return;
			this.assigned = assignments.assignments ?? [];
			const chosen = this.classes.find( ( c ) => c.id === classId );
			const name = chosen?.name ?? 'this class';
			await this.join.show( chosen ?? null );
			if ( load !== this.loads ) return;
			this.childrenNote.textContent = kids.length ? `In the class: ${ kids.map( ( kid ) => kid.display_name ).join( ', ' ) }.` : 'No children in this class yet.';
			this.assignedNote.textContent = this.assigned.length > 0 ? `${ name } has this lesson.` : `${ name } does not have this lesson yet.`;
			this.assignButton.disabled = this.assigned.length > 0;
			this.show( practiceRows( lists.flatMap( ( list ) => list.records ?? [] ), kids, lesson.items ) );

		} catch ( error ) {

			if ( load === this.loads ) this.showError( `The practice could not be loaded: ${ error.message }` );

		}

	}

	async assign() {

		const classId = this.classId;
		if ( ! this.lesson || classId === null ) return;
		this.assignButton.disabled = true;
		try {

			await this.api.post( 'assignments', { lesson_id: this.lesson.id, class_id: classId } );

		} catch ( error ) {

			this.assignButton.disabled = false;
			this.showError( `The lesson could not be assigned: ${ error.message }` );
			return;

		}

		await this.refresh();

	}

	show( rows ) {

		this.rows = rows;
		this.table.replaceChildren( ...rows.map( ( row ) => h( 'li', { className: 'lr-record' },
			picture( row.child.avatar, { label: row.child.avatar } ),
			h( 'span', { className: 'lr-record-name' }, row.child.display_name ),
			h( 'span', { className: 'lr-record-target' }, row.target ),
			row.rating ? picture( row.rating.face, { label: `${ row.rating.label } (${ row.ratedBy })`, className: 'cp-picture lr-face' } ) : h( 'span', { className: 'lr-face' }, '–' ),
			h( 'span', { className: 'lr-record-when' }, `${ shortTime( row.when ) }${ row.replays ? `, ${ row.replays } replay${ row.replays === 1 ? '' : 's' }` : '' }` ),
		) ) );
		if ( rows.length === 0 ) this.table.append( h( 'li', { className: 'lr-note' }, 'No practice of this lesson yet.' ) );

	}

	showError( message ) {

		this.error.textContent = message;
		this.error.hidden = ! message;

	}

	/** What window.glasshead.runner.panel reports. */
	report() {

		return {
			classId: this.classId, classes: this.classes.map( ( c ) => c.name ), assigned: this.assigned.length > 0,
			records: this.rows.map( ( row ) => ( { id: row.id, child: row.child.display_name, item: row.item, rating: row.rating?.rating ?? null, replays: row.replays } ) ),
			sharing: this.sharing.report(), join: this.join.report(),
		};

	}

}
