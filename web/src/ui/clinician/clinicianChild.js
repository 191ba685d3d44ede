// A child's history in the clinician view: choose a child of the caseload (the classes the
// clinician owns, GET /classes and GET /children), see every go they had at a lesson item
// (GET /practice?child_id=, newest first, with the item's target from the lesson) and their EPG
// recordings (GET /epg/recordings?child_id=), open a recording beside the target, and export the
// practice as CSV (GET /children/{id}/practice.csv) and a recording in the formats the server
// exports (GET /epg/recordings/{id}/export). The goes the child said into the microphone are
// plotted over the sessions (AttemptPlot.js), and the table says what each one measured, with a
// player for each go whose sound was kept (AttemptSound.js). The switch that keeps the sound of the
// child's goes is at the top (RecordingSwitch.js). The pure parts (the choices, the rows, the
// series, the switch in words) are in clinicianChildRows.js.

import { api as pageApi } from '../../api.js';
import { h } from '../shared/dom.js';
import { childChoices, EXPORT_FORMATS, measuredSeries, practiceRows, recordingExportPath } from './clinicianChildRows.js';
import { AttemptPlot } from './AttemptPlot.js';
import { AttemptSound } from './AttemptSound.js';
import { RecordingSwitch } from './RecordingSwitch.js';
import { downloadFile } from '../shared/download.js';
import './clinicianChild.css';

export class ChildHistory {

	/**
	 * @param {{ api?: object, onOpen?: ( id: number ) => void, download?: Function }} options
	 *   `onOpen( recordingId )` shows a recording in the view; `download( path, name )` saves a file
	 */
	constructor( { api = pageApi, onOpen = () => {}, download = downloadFile } = {} ) {

		this.api = api;
		this.onOpen = onOpen;
		this.download = download;
		this.lessons = new Map();
		this.state = { loaded: false, child: null, practice: 0, measured: 0, recordings: [], error: null };
		this.select = h( 'select', { 'aria-label': 'Child', className: 'cc-select', onChange: () => this.choose( this.select.value ) } );
		this.csvButton = h( 'button', { type: 'button', disabled: '', onClick: () => this.exportCsv() }, 'Export practice (CSV)' );
		this.status = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' }, 'Loading your caseload…' );
		this.table = h( 'table', { className: 'cv-table cc-practice', 'aria-label': 'Practice history' } );
		this.recordings = h( 'ul', { className: 'cc-recordings', 'aria-label': 'Recordings of the child' } );
		this.attempts = new AttemptPlot();
		this.recordingSwitch = new RecordingSwitch( { api } );
		this.sound = new AttemptSound( { api } );
		this.element = h( 'figure', { className: 'cv-card cc-child', 'aria-label': 'A child’s history' },
			h( 'figcaption', {}, 'A child’s history' ),
			h( 'div', { className: 'cc-bar' }, h( 'label', {}, 'Child ', this.select ), this.csvButton ),
			this.status, this.recordingSwitch.element,
			h( 'h3', { className: 'cc-heading' }, 'Practice' ), this.table,
			h( 'h3', { className: 'cc-heading' }, 'Spoken goes' ), this.attempts.element,
			h( 'h3', { className: 'cc-heading' }, 'Recordings' ), this.recordings );

	}

	/** What window.glasshead.clinician.child reports. */
	report() {

		return { ...this.state, options: [ ...this.select.options ].map( ( o ) => o.value ).filter( Boolean ), recording: this.recordingSwitch.report(), sound: this.sound.report() };

	}

	/** List the children of the caseload. */
	async load() {

		try {

			const [ classes, children ] = await Promise.all( [ this.api.get( 'classes?limit=1000' ), this.api.get( 'children?limit=1000' ) ] );
			const groups = childChoices( classes.classes, children.children );
			this.select.replaceChildren( h( 'option', { value: '' }, groups.length ? 'Choose a child' : 'No children in your caseload' ),
				...groups.map( ( group ) => h( 'optgroup', { label: group.label }, ...group.children.map( ( c ) => h( 'option', { value: c.value }, c.label ) ) ) ) );
			this.say( groups.length ? '' : 'Make a caseload and add children to it to follow them here.' );
			this.state.loaded = true;

		} catch ( error ) {

			this.fail( error );

		}

	}

	/** Show child `value` (an id as a string; '' for none). */
	async choose( value ) {

		const id = value ? Number( value ) : null;
		this.state = { ...this.state, child: id, practice: 0, recordings: [], error: null };
		this.csvButton.disabled = id === null;
		this.table.replaceChildren();
		this.recordings.replaceChildren();
		this.sound.dispose();
		this.recordingSwitch.load( id );
		if ( id === null ) return;
		this.say( 'Loading the child’s history…' );
		try {

			const [ practice, recordings ] = await Promise.all( [
				this.api.get( `practice?child_id=${ id }&limit=1000` ),
				this.api.get( `epg/recordings?child_id=${ id }&limit=1000` ),
			] );
			await this.loadLessons( practice.records );
			if ( this.state.child !== id ) return; // another child was chosen meanwhile
			this.showPractice( practiceRows( practice.records, this.lessons ), practice.total );
			this.state.measured = this.attempts.draw( measuredSeries( practice.records ) );
			this.showRecordings( recordings.recordings );
			this.say( '' );

		} catch ( error ) {

			if ( this.state.child === id ) this.fail( error );

		}

	}

	async loadLessons( records ) {

		const missing = [ ...new Set( records.map( ( r ) => r.lesson_id ) ) ].filter( ( id ) => ! this.lessons.has( id ) );
		const lessons = await Promise.all( missing.map( ( id ) => this.api.get( `lessons/${ id }` ).catch( () => null ) ) );
		missing.forEach( ( id, k ) => this.lessons.set( id, lessons[ k ] ) );

	}

	showPractice( rows, total ) {

		this.state.practice = total;
		const head = h( 'tr', {}, ...[ 'When (UTC)', 'Lesson', 'Item', 'Target', 'Replays', 'Rating', 'Heard' ].map( ( t ) => h( 'th', { scope: 'col' }, t ) ) );
		const body = rows.map( ( row ) => h( 'tr', { 'data-practice': String( row.id ) },
			...[ row.when, row.lesson, String( row.item ), row.target, String( row.replays ), row.rating ].map( ( t ) => h( 'td', {}, t ) ),
			h( 'td', {}, h( 'span', { className: 'cc-heard' }, ...( row.heard ? [ h( 'span', {}, row.heard ) ] : [] ), ...( row.audio ? [ this.sound.button( row.id, row.when ) ] : [] ) ) ) ) );
		this.table.replaceChildren( h( 'thead', {}, head ), h( 'tbody', {}, ...( body.length ? body : [ h( 'tr', {}, h( 'td', { colspan: '7' }, 'No practice yet.' ) ) ] ) ) );

	}

	showRecordings( recordings ) {

		this.state.recordings = recordings.map( ( r ) => r.id );
		const item = ( r ) => h( 'li', {},
			h( 'span', { className: 'cc-name', title: r.name }, `${ r.name }: ${ r.n_frames } frames, ${ r.duration_s.toFixed( 2 ) } s` ),
			h( 'button', { type: 'button', onClick: () => this.onOpen( r.id ) }, 'Compare' ),
			...EXPORT_FORMATS.map( ( f ) => h( 'button', {
				type: 'button', 'aria-label': `Export ${ r.name } as ${ f.label }`, onClick: () => this.exportRecording( r, f.format ),
			}, f.label ) ) );
		this.recordings.replaceChildren( ...( recordings.length ? recordings.map( item ) : [ h( 'li', {}, 'No recordings yet: import one above for this child.' ) ] ) );

	}

	async exportCsv() {

		const id = this.state.child;
		if ( id === null ) return;
		await this.save( `children/${ id }/practice.csv`, `child-${ id }-practice.csv` );

	}

	async exportRecording( recording, format ) {

		await this.save( recordingExportPath( recording.id, format ), `recording-${ recording.id }` );

	}

	async save( path, fallback ) {

		try {

			const name = await this.download( path, fallback );
			this.say( `Saved ${ name }.` );

		} catch ( error ) {

			this.fail( error );

		}

	}

	/** Let go of the sounds opened (the view is leaving). */
	dispose() {

		this.sound.dispose();

	}

	say( text ) {

		this.status.textContent = text;

	}

	fail( error ) {

		this.state.error = error.message;
		this.say( error.message );

	}

}
